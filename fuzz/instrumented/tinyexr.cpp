// tinyexr's implementation, compiled from Debian's own header (libtinyexr-dev,
// the same version as the shared library the normal build links) into
// wavepath_image in sanitizer and fuzz builds, with their flags
// (cmake/InstrumentedDeps.cmake says why). Settings as in Debian's build:
// zlib for ZIP, PIZ on, no threads.
#define TINYEXR_IMPLEMENTATION
#define TINYEXR_USE_MINIZ 0
#include <zlib.h>

#include <tinyexr.h>
