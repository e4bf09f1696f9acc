#!/usr/bin/env python3
"""Two closed rooms side by side, a lamp in A only and no opening between them: every watt in B is a leak.

closed_rooms_obj.py OUT.obj THICKNESS [SHIFT]   THICKNESS of the shared wall (0: coincident faces); SHIFT
slides B along the wall, so that each room's side wall meets the other's wall mid-span. Cells A and B
are `g cell:` groups, so `cpgi compare-light` reports each (bench/RESULTS.md, "Light through a
zero-thickness wall on the GL engine")."""
import sys
out, t = sys.argv[1], float(sys.argv[2])
shift = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
V, F = [], []
def quad(p0, p1, p2, p3, n, mat):
    # wind so that (p1-p0)x(p2-p0) points along n
    a = [p1[i]-p0[i] for i in range(3)]; b = [p2[i]-p0[i] for i in range(3)]
    c = [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
    pts = [p0, p1, p2, p3] if sum(c[i]*n[i] for i in range(3)) > 0 else [p3, p2, p1, p0]
    base = len(V) + 1
    V.extend(pts); F.append((mat, [base, base+1, base+2, base+3]))
def room(x0, x1, z0, z1, h, mat, name):
    F.append(("group", name))
    quad((x0,0,z0),(x1,0,z0),(x1,0,z1),(x0,0,z1),(0,1,0),mat)      # floor
    quad((x0,h,z0),(x1,h,z0),(x1,h,z1),(x0,h,z1),(0,-1,0),mat)     # ceiling
    quad((x0,0,z0),(x0,h,z0),(x0,h,z1),(x0,0,z1),(1,0,0),mat)      # -x wall
    quad((x1,0,z0),(x1,h,z0),(x1,h,z1),(x1,0,z1),(-1,0,0),mat)     # +x wall
    quad((x0,0,z0),(x1,0,z0),(x1,h,z0),(x0,h,z0),(0,0,1),mat)      # -z wall
    quad((x0,0,z1),(x1,0,z1),(x1,h,z1),(x0,h,z1),(0,0,-1),mat)     # +z wall
h = 2.6
room(-4, 0, 0, 4, h, "white", "A")
room(t, 4 + t, shift, 4 + shift, h, "white", "B")
F.append(("group","A"))
quad((-2.5,h-0.01,1.5),(-1.5,h-0.01,1.5),(-1.5,h-0.01,2.5),(-2.5,h-0.01,2.5),(0,-1,0),"light")
with open(out.replace('.obj','.mtl'),'w') as m:
    m.write("newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.8 0.8 0.8\nKe 100 100 100\n")
with open(out,'w') as o:
    o.write("mtllib %s\n" % out.split('/')[-1].replace('.obj','.mtl'))
    for v in V: o.write("v %g %g %g\n" % v)
    cur = None
    for mat, f in F:
        if mat == "group": o.write("g cell:%s\n" % f); continue
        if mat != cur: o.write("usemtl %s\n" % mat); cur = mat
        o.write("f %s\n" % " ".join(map(str, f)))
