#!/usr/bin/env python3
"""Two closed rooms side by side, a lamp in A only and no opening between them: every watt in B is a leak.

closed_rooms_obj.py OUT.obj THICKNESS [SHIFT]   THICKNESS of the shared wall (0: coincident faces); SHIFT
slides B along the wall, so that each room's side wall meets the other's wall mid-span. Cells A and B
are `g cell:` groups, so `cpgi compare-light` reports each (bench/RESULTS.md, "Light through a
zero-thickness wall on the GL engine")."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cell_obj import CellObj  # noqa: E402

out, t = sys.argv[1], float(sys.argv[2])
shift = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
obj = CellObj()
quad = obj.quad
def room(x0, x1, z0, z1, h, mat, name):
    obj.group(name)
    quad((x0,0,z0),(x1,0,z0),(x1,0,z1),(x0,0,z1),(0,1,0),mat)      # floor
    quad((x0,h,z0),(x1,h,z0),(x1,h,z1),(x0,h,z1),(0,-1,0),mat)     # ceiling
    quad((x0,0,z0),(x0,h,z0),(x0,h,z1),(x0,0,z1),(1,0,0),mat)      # -x wall
    quad((x1,0,z0),(x1,h,z0),(x1,h,z1),(x1,0,z1),(-1,0,0),mat)     # +x wall
    quad((x0,0,z0),(x1,0,z0),(x1,h,z0),(x0,h,z0),(0,0,1),mat)      # -z wall
    quad((x0,0,z1),(x1,0,z1),(x1,h,z1),(x0,h,z1),(0,0,-1),mat)     # +z wall
h = 2.6
room(-4, 0, 0, 4, h, "white", "A")
room(t, 4 + t, shift, 4 + shift, h, "white", "B")
obj.group("A")
quad((-2.5,h-0.01,1.5),(-1.5,h-0.01,1.5),(-1.5,h-0.01,2.5),(-2.5,h-0.01,2.5),(0,-1,0),"light")
obj.write(out, "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.8 0.8 0.8\nKe 100 100 100\n")
