#!/usr/bin/env python3
# Where a converted Quake III level is open (issue 46): the OBJ's triangles marked into voxels of VOXEL
# metres (points every third of a voxel), a 6-connected flood of the empty voxels from the grid's border,
# then for each spawn point of the BSP (info_player_*, team_CTF_*) whether the flood reaches it, and the
# path from the first one reached back to the border: the hole, as q3map2's .lin file shows a leak. A
# level the decomposition takes for the outside is open this way (bench/RESULTS.md, "Eight OpenArena
# 0.8.5/0.8.8 maps"). Pure Python, a few seconds at 1 m on a 4 000-triangle map; OBJ from q3bsp_to_obj at
# its default 0.03 m a unit.
#   bench/q3_leak_path.py MAP.obj MAP.bsp VOXEL
import sys,math,collections,struct,re
obj,bsp,h=sys.argv[1],sys.argv[2],float(sys.argv[3])
V=[];T=[]
for l in open(obj):
    if l.startswith('v '): V.append(tuple(float(x) for x in l.split()[1:4]))
    elif l.startswith('f '): T.append([int(x.split('/')[0])-1 for x in l.split()[1:]])
lo=[min(v[k] for v in V)-2*h for k in range(3)]; hi=[max(v[k] for v in V)+2*h for k in range(3)]
n=[int(math.ceil((hi[k]-lo[k])/h)) for k in range(3)]
solid=bytearray(n[0]*n[1]*n[2])
def idx(i,j,k): return (i*n[1]+j)*n[2]+k
def mark(p):
    i,j,k=(int((p[d]-lo[d])/h) for d in range(3))
    solid[idx(i,j,k)]=1
step=h/3
for t in T:
    a,b,c=(V[i] for i in t[:3])
    e1=[b[d]-a[d] for d in range(3)]; e2=[c[d]-a[d] for d in range(3)]
    m=max(1,int(math.ceil(max(math.dist(a,b),math.dist(a,c),math.dist(b,c))/step)))
    for u in range(m+1):
        for v in range(m+1-u):
            mark([a[d]+e1[d]*u/m+e2[d]*v/m for d in range(3)])
par={}
q=collections.deque()
for i in range(n[0]):
    for j in range(n[1]):
        for k in range(n[2]):
            if i in (0,n[0]-1) or j in (0,n[1]-1) or k in (0,n[2]-1):
                x=idx(i,j,k)
                if not solid[x]: par[x]=-1; q.append((i,j,k))
while q:
    i,j,k=q.popleft()
    for di,dj,dk in ((1,0,0),(-1,0,0),(0,1,0),(0,-1,0),(0,0,1),(0,0,-1)):
        a,b,c=i+di,j+dj,k+dk
        if 0<=a<n[0] and 0<=b<n[1] and 0<=c<n[2]:
            x=idx(a,b,c)
            if x not in par and not solid[x]: par[x]=idx(i,j,k); q.append((a,b,c))
data=open(bsp,'rb').read(); off,ln=struct.unpack_from('<ii',data,8); ents=data[off:off+ln].decode('latin1')
spawns=[]
for e in re.findall(r'\{[^{}]*\}',ents):
    c=re.search(r'"classname"\s+"([^"]+)"',e); o=re.search(r'"origin"\s+"([^"]+)"',e)
    if c and o and c.group(1).startswith(('info_player','team_CTF')):
        x,y,z=map(float,o.group(1).split()); spawns.append((c.group(1),(x*0.03,z*0.03,-y*0.03)))
print('grid',n,'solid',sum(solid),'flooded',len(par))
def cen(x):
    k=x%n[2]; j=(x//n[2])%n[1]; i=x//(n[1]*n[2]); return tuple(round(lo[d]+(v+0.5)*h,1) for d,v in enumerate((i,j,k)))
first=None
for name,p in spawns:
    x=idx(*(int((p[d]-lo[d])/h) for d in range(3)))
    r=x in par; print(name,[round(c,1) for c in p],'reached from the border' if r else 'sealed')
    if r and first is None: first=x
if first is not None:
    path=[];x=first
    while x!=-1: path.append(cen(x)); x=par[x]
    print('path length',len(path)); print('last 25 voxels to the border:',path[-25:])
