# Content for the undecodable-texture test: the glTF corpus, written by its generator.
file(REMOVE_RECURSE ${OUT}/corpus)
execute_process(COMMAND ${CORPUS} ${OUT}/corpus RESULT_VARIABLE corpus_rc OUTPUT_QUIET)
if(NOT corpus_rc EQUAL 0)
  message(FATAL_ERROR "gltf_corpus ${OUT}/corpus: exit code ${corpus_rc}")
endif()
