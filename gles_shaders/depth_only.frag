// Depth prepass: only the depth buffer is written.
precision lowp float;
void main() {}
