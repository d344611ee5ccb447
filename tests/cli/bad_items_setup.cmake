# Content for the bad-items test: a missing scene, a corrupt .glb and a valid one, in one playlist.
set(dir ${OUT}/bad-items)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/corrupt.glb "glTF this is not")
file(COPY ${SHARED}/scenes/spot.glb DESTINATION ${dir})
file(WRITE ${dir}/list.toml "loop = true
fade = 0.0
[[item]]
scene = \"missing.glb\"
duration = 0.5
[[item]]
scene = \"corrupt.glb\"
duration = 0.5
[[item]]
scene = \"spot.glb\"
duration = 0.5
camera = { motion = \"turntable\", period = 20.0, elevation = 15.0, distance = 1.1 }
ao = { estimator = \"horizon\", samples = 32 }
")
