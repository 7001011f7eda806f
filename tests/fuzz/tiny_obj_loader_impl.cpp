// tinyobjloader's implementation, compiled into the fuzz targets with their instrumentation so that
// ASan, UBSan and libFuzzer's coverage see inside the parser too. The host links Debian's
// libtinyobjloader instead, which is built from this same header (libtinyobjloader-dev 2.0.0~rc10).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
