// Precision and helpers shared by the compute passes.
#ifdef AO_MEDIUMP
precision mediump float;
#else
precision highp float;
#endif
precision highp int;
precision highp sampler2D;
precision highp image2D;
