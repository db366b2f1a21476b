#version 330 core
// Mesh geometry stage: gives each corner its distances (in pixels) to the three edges of its
// triangle, so the fragment stage can draw a wireframe whose width is constant on screen at
// any zoom, in the same pass as the surface.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform vec2 u_viewport_size;

in VertexData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
  vec3 world_position;
} v_in[];

out FragmentData {
  vec3 view_position;
  vec3 view_normal;
  float scalar;
  vec3 world_position;
  noperspective vec3 edge_distance;
  // Categorical fields (valence, level): the three corners' values and where in the
  // triangle the fragment is, so it takes its nearest corner's value unblended.
  flat vec3 corner_scalars;
  vec3 barycentric;
} g_out;

vec2 to_pixels(vec4 clip) { return 0.5 * u_viewport_size * clip.xy / clip.w; }

void main() {
  vec2 p0 = to_pixels(gl_in[0].gl_Position);
  vec2 p1 = to_pixels(gl_in[1].gl_Position);
  vec2 p2 = to_pixels(gl_in[2].gl_Position);
  // Height of each corner above its opposite edge: twice the area over the edge's length.
  float area2 = abs((p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x));
  vec3 heights = area2 / max(vec3(length(p2 - p1), length(p2 - p0), length(p1 - p0)), 1e-6);
  // A corner behind the eye would give meaningless pixel positions: no wire then.
  if (gl_in[0].gl_Position.w <= 0.0 || gl_in[1].gl_Position.w <= 0.0 ||
      gl_in[2].gl_Position.w <= 0.0) {
    heights = vec3(1e6);
  }
  for (int i = 0; i < 3; ++i) {
    g_out.view_position = v_in[i].view_position;
    g_out.view_normal = v_in[i].view_normal;
    g_out.scalar = v_in[i].scalar;
    g_out.world_position = v_in[i].world_position;
    g_out.edge_distance = vec3(0.0);
    g_out.edge_distance[i] = heights[i];
    g_out.corner_scalars = vec3(v_in[0].scalar, v_in[1].scalar, v_in[2].scalar);
    g_out.barycentric = vec3(0.0);
    g_out.barycentric[i] = 1.0;
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
