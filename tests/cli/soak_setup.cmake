# The soak playlist with a shared scene beside it (a playlist's files stay inside its folder).
set(dir ${OUT}/soak)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(COPY ${SOURCE}/list.toml ${SHARED}/scenes/spot.glb DESTINATION ${dir})
