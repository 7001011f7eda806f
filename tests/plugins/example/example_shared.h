// The example's block, one declaration for example.cpp and example.glsl.
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(example)
SHADOWLAB_UNIFORM_BLOCK(ExampleUniforms, 2) { float uDarkness, uPad0, uPad1, uPad2; };
SHADOWLAB_SHARED_END
