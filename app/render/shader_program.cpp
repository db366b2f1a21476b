#include "app/render/shader_program.h"

#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "app/render/gl_api.h"
#include "app/render/shader_sources.h"

namespace dynamesh {
namespace {

GLuint compile_stage(GLenum stage, std::string_view file) {
  const std::string_view text = shader_source(file);
  if (text.empty()) throw std::runtime_error("shader file not embedded: " + std::string(file));
  const GLuint shader = gl::CreateShader(stage);
  const char* data = text.data();
  const GLint length = static_cast<GLint>(text.size());
  gl::ShaderSource(shader, 1, &data, &length);
  gl::CompileShader(shader);
  GLint ok = GL_FALSE;
  gl::GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::vector<char> log(4096);
    gl::GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl::DeleteShader(shader);
    throw std::runtime_error("cannot compile " + std::string(file) + ": " + log.data());
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(std::string_view vertex_file, std::string_view geometry_file,
                             std::string_view fragment_file) {
  std::vector<GLuint> stages{compile_stage(GL_VERTEX_SHADER, vertex_file),
                             compile_stage(GL_FRAGMENT_SHADER, fragment_file)};
  if (!geometry_file.empty()) stages.push_back(compile_stage(GL_GEOMETRY_SHADER, geometry_file));
  id_ = gl::CreateProgram();
  for (GLuint s : stages) gl::AttachShader(id_, s);
  gl::LinkProgram(id_);
  for (GLuint s : stages) gl::DeleteShader(s);  // flagged; freed with the program
  GLint ok = GL_FALSE;
  gl::GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::vector<char> log(4096);
    gl::GetProgramInfoLog(id_, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl::DeleteProgram(id_);
    throw std::runtime_error("cannot link " + std::string(vertex_file) + ": " + log.data());
  }
}

ShaderProgram::~ShaderProgram() {
  if (id_ != 0) gl::DeleteProgram(id_);
}

void ShaderProgram::use() const {
  gl::UseProgram(id_);
}

int ShaderProgram::location(const char* name) {
  auto it = locations_.find(name);
  if (it == locations_.end())
    it = locations_.emplace(name, gl::GetUniformLocation(id_, name)).first;
  return it->second;
}

void ShaderProgram::set(const char* name, int value) {
  gl::Uniform1i(location(name), value);
}
void ShaderProgram::set(const char* name, float value) {
  gl::Uniform1f(location(name), value);
}
void ShaderProgram::set(const char* name, const glm::vec2& v) {
  gl::Uniform2f(location(name), v.x, v.y);
}
void ShaderProgram::set(const char* name, const glm::vec3& v) {
  gl::Uniform3f(location(name), v.x, v.y, v.z);
}
void ShaderProgram::set(const char* name, const glm::mat3& m) {
  gl::UniformMatrix3fv(location(name), 1, GL_FALSE, glm::value_ptr(m));
}
void ShaderProgram::set(const char* name, const glm::mat4& m) {
  gl::UniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace dynamesh
