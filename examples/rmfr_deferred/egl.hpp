#pragma once
#include <string>
/// Makes a headless GL 4.5 core context current on this thread; "" or what failed.
std::string make_headless_gl_context();
