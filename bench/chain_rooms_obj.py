#!/usr/bin/env python3
"""A chain of N rooms along +x, 4 x 4 x 2.6 m, walls T thick (0: coincident faces), a door W wide in each
shared wall, centred or D from the side wall, a 1 m^2 lamp of 100 W/m^2 under R1's ceiling only; cells
R1..RN as `g cell:` groups (bench/RESULTS.md, "The dim rooms' bias apart").

  chain_rooms_obj.py OUT.obj [N] [T] [W] [D]"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cell_obj import CellObj  # noqa: E402

out = sys.argv[1]
N = int(sys.argv[2]) if len(sys.argv) > 2 else 4
T = float(sys.argv[3]) if len(sys.argv) > 3 else 0.2
W = float(sys.argv[4]) if len(sys.argv) > 4 else 1.0
D = float(sys.argv[5]) if len(sys.argv) > 5 else -1.0  # door start from the side wall; <0: centred
h, dh, L = 2.6, 2.1, 4.0
obj = CellObj()
quad = obj.quad
def doorSpan(z0, z1):
    if D < 0: zc = 0.5*(z0+z1); return zc-W/2, zc+W/2
    return z0+D, z0+D+W
def xwall(x, sgn, z0, z1, door, mat):
    """A wall perpendicular to x at x, facing sgn, over z0..z1, with a door centred if door."""
    n = (sgn, 0, 0)
    if not door:
        quad((x,0,z0),(x,h,z0),(x,h,z1),(x,0,z1),n,mat); return
    d0, d1 = doorSpan(z0, z1)
    quad((x,0,z0),(x,h,z0),(x,h,d0),(x,0,d0),n,mat)
    quad((x,0,d1),(x,h,d1),(x,h,z1),(x,0,z1),n,mat)
    quad((x,dh,d0),(x,h,d0),(x,h,d1),(x,dh,d1),n,mat)
for r in range(N):
    x0 = r*(L+T); x1 = x0+L; z0, z1 = 0.0, L
    obj.group("R%d" % (r+1))
    quad((x0,0,z0),(x1,0,z0),(x1,0,z1),(x0,0,z1),(0,1,0),"floor")
    quad((x0,h,z0),(x1,h,z0),(x1,h,z1),(x0,h,z1),(0,-1,0),"ceiling")
    xwall(x0, 1, z0, z1, r > 0, "wall")
    xwall(x1, -1, z0, z1, r < N-1, "wall")
    quad((x0,0,z0),(x1,0,z0),(x1,h,z0),(x0,h,z0),(0,0,1),"wall")
    quad((x0,0,z1),(x1,0,z1),(x1,h,z1),(x0,h,z1),(0,0,-1),"wall")
    if r == 0:
        c = 0.5*L
        quad((x0+c-.5,h-.01,c-.5),(x0+c+.5,h-.01,c-.5),(x0+c+.5,h-.01,c+.5),(x0+c-.5,h-.01,c+.5),(0,-1,0),"light")
    if r < N-1 and T > 0:  # the door's reveal, given to the room on its low side
        a, b = x1, x1+T; d0, d1 = doorSpan(0.0, L)
        quad((a,0,d0),(b,0,d0),(b,dh,d0),(a,dh,d0),(0,0,1),"reveal")
        quad((a,0,d1),(b,0,d1),(b,dh,d1),(a,dh,d1),(0,0,-1),"reveal")
        quad((a,dh,d0),(b,dh,d0),(b,dh,d1),(a,dh,d1),(0,-1,0),"reveal")
        quad((a,0,d0),(b,0,d0),(b,0,d1),(a,0,d1),(0,1,0),"floor")
obj.write(out, "newmtl wall\nKd 0.7 0.7 0.7\nnewmtl floor\nKd 0.5 0.5 0.5\nnewmtl ceiling\nKd 0.8 0.8 0.8\n"
            "newmtl reveal\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.8 0.8 0.8\nKe 100 100 100\n")
