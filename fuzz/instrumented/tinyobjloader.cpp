// tinyobjloader's implementation, compiled from Debian's own header
// (libtinyobjloader-dev, the same version as libtinyobjloader_double.so, which
// the normal build links) into wavepath_scene in sanitizer and fuzz builds,
// with their flags (cmake/InstrumentedDeps.cmake says why).
// TINYOBJLOADER_USE_DOUBLE comes from the tinyobjloader::tinyobjloader_double
// target, as for the shared library.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
