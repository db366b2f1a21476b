// A linked GLSL program built from embedded shader files, with uniform setters that look
// locations up by name (programs here are small; lookups are cached).
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>

#include <glm/glm.hpp>

namespace dynamesh {

class ShaderProgram {
 public:
  // Compiles and links the named files of shaders/ (geometry may be empty). Throws
  // std::runtime_error with the compiler's log when a stage does not compile or link.
  ShaderProgram(std::string_view vertex_file, std::string_view geometry_file,
                std::string_view fragment_file);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const;
  void set(const char* name, int value);
  void set(const char* name, bool value) { set(name, value ? 1 : 0); }
  void set(const char* name, float value);
  void set(const char* name, const glm::vec2& value);
  void set(const char* name, const glm::vec3& value);
  void set(const char* name, const glm::mat3& value);
  void set(const char* name, const glm::mat4& value);

 private:
  int location(const char* name);

  unsigned id_ = 0;
  std::unordered_map<std::string, int> locations_;
};

}  // namespace dynamesh
