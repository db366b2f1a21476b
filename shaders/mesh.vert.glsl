#version 330 core
// Mesh vertex stage: to view space; the scalar of the active colour mode and the world
// position (where a volume is sampled, per fragment) ride along.
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
  vec3 world_position;
} v_out;

void main() {
  vec4 view = u_model_view * vec4(a_position, 1.0);
  v_out.view_position = view.xyz;
  v_out.view_normal = u_normal_matrix * a_normal;
  v_out.scalar = a_scalar;
  v_out.world_position = a_position;
  gl_Position = u_projection * view;
}
