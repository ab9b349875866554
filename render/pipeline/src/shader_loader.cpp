#include "foveal/render/shader_loader.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

#include "foveal/core/data_paths.hpp"
#include "foveal/rmfr.hpp"

namespace foveal::gl {

namespace {

constexpr int kMaxIncludeDepth = 16;

Result<std::string> read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return io_error(path + ": cannot open shader file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Expands `path` into `out`, giving each file a source-string number.
Status expand_into(const std::string& root, const std::string& path, int depth, std::vector<std::string>& files,
                   std::string& out, const std::vector<VirtualFile>& virtual_files) {
  if (depth > kMaxIncludeDepth) return bad_input(path + ": #include nested deeper than 16 (a cycle?)");
  // foveal-rmfr's GLSL (`foveal/...`) comes from the library itself: one copy of RMFR's
  // mapping for the compositor's shaders and the library's passes.
  const std::string_view builtin = rmfr::glsl_file(path);
  std::string name = builtin.empty() ? root + "/" + path : "foveal-rmfr:" + path;
  auto text = builtin.empty() ? Result<std::string>(std::string()) : Result<std::string>(std::string(builtin));
  if (path.rfind("method/", 0) == 0) {  // the caller's, or empty
    name = path;
    for (const VirtualFile& v : virtual_files)
      if (v.name == path) text = v.text;
  } else if (builtin.empty()) {
    text = read_text(name);
  }
  if (!text) return text.error();
  const int index = static_cast<int>(files.size());
  files.push_back(name);
  out += "#line 1 " + std::to_string(index) + "\n";
  std::istringstream lines(*text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::size_t p = line.find_first_not_of(" \t");
    if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
      const std::size_t a = line.find('"', p), b = a == std::string::npos ? a : line.find('"', a + 1);
      if (b == std::string::npos)
        return bad_input(root + "/" + path + ":" + std::to_string(number) + ": expected #include \"file\"");
      if (Status s = expand_into(root, line.substr(a + 1, b - a - 1), depth + 1, files, out, virtual_files); !s) return s;
      out += "#line " + std::to_string(number + 1) + " " + std::to_string(index) + "\n";
      continue;
    }
    out += line;
    out += '\n';
  }
  return {};
}

std::string shader_log(GLuint shader) {
  GLint len = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
  glGetShaderInfoLog(shader, len, nullptr, log.data());
  return log.c_str();
}

std::string program_log(GLuint program) {
  GLint len = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
  glGetProgramInfoLog(program, len, nullptr, log.data());
  return log.c_str();
}

// Parses an unsigned integer at s[i], advancing i; -1 if none.
long parse_uint(const std::string& s, std::size_t& i) {
  if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) return -1;
  long v = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])) && v < 1000000) v = v * 10 + (s[i++] - '0');
  return v;
}

}  // namespace

std::string map_info_log(const std::string& log, const std::vector<std::string>& files) {
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    std::size_t i = 0;
    const long src = parse_uint(line, i);
    long number = -1;
    std::size_t rest = 0;
    if (src >= 0 && i < line.size() && line[i] == ':') {  // Mesa: 0:12(5): msg
      ++i;
      number = parse_uint(line, i);
      if (number >= 0 && i < line.size() && line[i] == '(') {
        rest = line.find("):", i);
        rest = rest == std::string::npos ? 0 : rest + 2;
      } else {
        number = -1;
      }
    } else if (src >= 0 && i < line.size() && line[i] == '(') {  // NVIDIA: 0(12) : msg
      ++i;
      number = parse_uint(line, i);
      rest = line.find(':', i);
      rest = rest == std::string::npos ? 0 : rest + 1;
    }
    if (number >= 0 && rest > 0 && static_cast<std::size_t>(src) < files.size()) {
      std::size_t m = line.find_first_not_of(' ', rest);
      out += files[static_cast<std::size_t>(src)] + ":" + std::to_string(number) + ": " +
             line.substr(m == std::string::npos ? line.size() : m) + "\n";
    } else if (!line.empty()) {
      out += line + "\n";
    }
  }
  return out;
}

ShaderLoader::ShaderLoader(std::string root) : root_(root.empty() ? data_path("shaders") : std::move(root)) {}

Result<std::string> ShaderLoader::expand(const std::string& path, std::vector<std::string>& files,
                                         const std::vector<VirtualFile>& virtual_files) const {
  std::string out;
  if (Status s = expand_into(root_, path, 0, files, out, virtual_files); !s) return s.error();
  return out;
}

Result<Program> ShaderLoader::program(const std::vector<ShaderStage>& stages, const std::string& defines,
                                      const std::vector<VirtualFile>& virtual_files) const {
  Program program = Program::create();
  std::vector<Shader> shaders;
  std::string names;
  for (const ShaderStage& stage : stages) {
    std::vector<std::string> files;
    auto body = expand(stage.path, files, virtual_files);
    if (!body) return body.error();
    const std::string source = "#version 450 core\n" + defines + *body;
    Shader shader(glCreateShader(stage.type));
    const char* text = source.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) return bad_input("shader compile error:\n" + map_info_log(shader_log(shader.id()), files));
    glAttachShader(program.id(), shader.id());
    names += (names.empty() ? "" : " + ") + root_ + "/" + stage.path;
    shaders.push_back(std::move(shader));
  }
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) return bad_input(names + ": shader link error:\n" + program_log(program.id()));
  for (const Shader& s : shaders) glDetachShader(program.id(), s.id());
  return program;
}

}  // namespace foveal::gl
