// Planar shadows: the flattened caster marks its pixels as shadowed.
layout(location = 0) out float outMask;

void main() {
    outMask = 0.0;
}
