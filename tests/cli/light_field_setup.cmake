# Content for the light field play test: a scene on a quilt display, one on optical modules, and one on
# a display file with an error (that item is skipped and reported; the others play).
set(dir ${OUT}/light-field)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/visual.json "{\"pitch\": {\"value\": 50}, \"slope\": {\"value\": -5}, \"center\": {\"value\": 0.1}, \"DPI\": {\"value\": 300},
 \"screenW\": {\"value\": 96}, \"screenH\": {\"value\": 128}, \"invView\": {\"value\": 1}}")
file(WRITE ${dir}/quilt.toml "type = \"quilt\"
calibration = \"visual.json\"
quilt = \"4x3\"
view_size = \"24x32\"
")
file(WRITE ${dir}/modules.toml "type = \"modules\"
[screen]
width = 1.6
height = 0.9
[observer]
distance = 2.5
[modules]
count = 4
x_first = -1.0
x_last = 1.0
z = -1.2
resolution = \"48x27\"
")
file(WRITE ${dir}/broken.toml "type = \"modules\"
[screen]
width = 1.6
height = 0.9
[observer]
distance = 2.5
[modules]
count = 0
")
file(WRITE ${dir}/list.toml "loop = true
fade = 0.0
[[item]]
scene = \"builtin:corner\"
duration = 1.0
display = \"quilt.toml\"
[[item]]
scene = \"builtin:spheres\"
duration = 1.0
display = \"modules.toml\"
[[item]]
scene = \"builtin:corner\"
duration = 1.0
display = \"broken.toml\"
")
