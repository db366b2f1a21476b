#version 330 core
// Mesh vertex stage: to view space; the scalar of the active colour mode rides along.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_scalar;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out VertexData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
} v_out;

void main() {
  vec4 view = u_model_view * vec4(a_position, 1.0);
  v_out.view_position = view.xyz;
  v_out.view_normal = u_normal_matrix * a_normal;
  v_out.scalar = a_scalar;
  gl_Position = u_projection * view;
}
