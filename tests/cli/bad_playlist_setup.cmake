set(dir ${OUT}/bad-playlist)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/list.toml "[[item]]
scene = \"builtin:demo\"
duration = \"long\"
")
