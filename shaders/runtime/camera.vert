#version 450
// The camera-in draw's full-screen triangle (three vertices, no vertex buffer): covers the viewport once.
void main() {
    const vec2 corner = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
