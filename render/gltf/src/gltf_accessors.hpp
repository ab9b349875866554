#pragma once
// A glTF accessor's elements, read with every byte checked before its output is
// allocated: the accessor's type and component type against what the use accepts, its
// elements inside its buffer view, the view inside its buffer (64-bit, no wrap), the
// output counted against the loader's decode budget. Messages: "FILE: PATH: what".
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "gltf_internal.hpp"

namespace foveal::render::detail {

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& m, std::string file, const GltfLimits& limits, DecodeBudget& budget)
      : m_(m), file_(std::move(file)), limits_(limits), budget_(budget) {}

  /// bad_input "FILE: PATH: what".
  Error fail(const std::string& path, const std::string& what) const { return bad_input(file_ + ": " + path + ": " + what); }

  /// Accessor `index` as n floats per element (normalised integers scaled as the spec
  /// says; no buffer view: all zeros), its component type one of `types`, each finite.
  Result<std::vector<float>> floats(int index, int n, std::initializer_list<int> types, const std::string& use);

  /// Index accessor `index` (unsigned byte, short or int, with a buffer view) as 32 bits.
  Result<std::vector<std::uint32_t>> indices(int index, const std::string& use);

 private:
  // Where an accessor's elements are: element i starts at base + stride * i.
  struct Span {
    const unsigned char* base = nullptr;  // null: no buffer view, all zeros
    std::size_t stride = 0, count = 0;
    int component_type = 0, comps = 0;
    bool normalized = false;
  };
  Result<Span> span(int index, int type, std::initializer_list<int> types, const std::string& use) const;

  const tinygltf::Model& m_;
  std::string file_;
  const GltfLimits& limits_;
  DecodeBudget& budget_;
};

}  // namespace foveal::render::detail
