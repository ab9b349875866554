// Fuzz builds only (FOVEAL_FUZZ): tinygltf 2.7 and stb_image compiled from Debian's
// headers into foveal::gltf, so ASan and UBSan see inside them as well. The normal
// build links Debian's shared libraries, which are not instrumented.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
