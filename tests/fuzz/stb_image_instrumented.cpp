// In the fuzz build, stb_image is compiled here from Debian's header so that
// libFuzzer sees its branches (Debian's libstb is not instrumented). The
// program's own definitions take precedence over the shared library's.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
