#version 450
// Per-primitive layer selection, as the multi-resolution caustic map does (Wyman 2008 Sec. 3.3).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) flat in int v_instance[];
layout(location = 0) flat out int g_layer;
void main() {
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gl_Layer = v_instance[0];
        g_layer = v_instance[0];
        EmitVertex();
    }
    EndPrimitive();
}
