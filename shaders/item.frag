flat in int vPatch;
layout(location = 0) out int outPatch;
void main() { outPatch = vPatch; }
