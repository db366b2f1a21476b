#version 330 core
// Mesh vertex stage straight into the fragment stage, for drawing without the wireframe:
// no geometry stage, which software renderers (llvmpipe) run slowly on one thread.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_scalar;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out FragmentData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
  noperspective vec3 edge_distance;
} v_out;

void main() {
  vec4 view = u_model_view * vec4(a_position, 1.0);
  v_out.view_position = view.xyz;
  v_out.view_normal = u_normal_matrix * a_normal;
  v_out.scalar = a_scalar;
  v_out.edge_distance = vec3(1e6);  // far from every edge: no wire
  gl_Position = u_projection * view;
}
