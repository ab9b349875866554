#pragma once
// GLSL programs from the files in shaders/, read at run time. Files hold no #version
// line (the loader adds "#version 450 core" and the caller's defines); a line
// `#include "path"` pulls in another file relative to the shader root (`foveal/...`
// names foveal-rmfr's GLSL, which comes from the library: foveal::rmfr::glsl_file; that
// is why the loader stands on the pipeline's floor, above foveal-rmfr, and not in
// render/gl). Compile and link errors are reported as "file:line: message" for the file
// the line came from. `method/...` names are virtual files the caller gives with the
// program (a described foveation method's kernel, foveal/image/method_description.hpp);
// one not given is empty.
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/render/gl_objects.hpp"

namespace foveal::gl {

struct ShaderStage {
  GLenum type;       ///< GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
  std::string path;  ///< relative to the shader root
};

/// Text an `#include "method/NAME"` line takes instead of a file.
struct VirtualFile {
  std::string name;  ///< "method/NAME"
  std::string text;
};

class ShaderLoader {
 public:
  /// `root` holds the shader files; default: data_path("shaders").
  explicit ShaderLoader(std::string root = {});

  /// Compiles and links. `defines` are inserted after #version (e.g. "#define X 1\n").
  /// Errors: a missing file (io, names it), a compile or link error (bad_input, with
  /// file:line of every message). Needs a current context.
  Result<Program> program(const std::vector<ShaderStage>& stages, const std::string& defines = {},
                          const std::vector<VirtualFile>& virtual_files = {}) const;

  /// The expanded source of one file with #line markers, and the file of each source
  /// number (index = GLSL source-string number). For tests and error mapping.
  Result<std::string> expand(const std::string& path, std::vector<std::string>& files,
                             const std::vector<VirtualFile>& virtual_files = {}) const;

  const std::string& root() const { return root_; }

 private:
  std::string root_;
};

/// Rewrites a driver's info log ("0:12(5): error..." from Mesa, "0(12) : error..." from
/// NVIDIA) so each message names files[N]:LINE. Lines it does not recognise stay as they are.
std::string map_info_log(const std::string& log, const std::vector<std::string>& files);

}  // namespace foveal::gl
