"""An OBJ of quads in `g cell:NAME` groups, with its .mtl beside it, for the bench's hand-made scenes
(chain_rooms_obj.py, closed_rooms_obj.py): cpgi reads each group as a cell."""


class CellObj:
    def __init__(self):
        self.vertices, self.faces = [], []  # faces: (material, [1-based indices]) or ("group", name)

    def group(self, name):
        self.faces.append(("group", name))

    def quad(self, p0, p1, p2, p3, n, mat):
        """The quad p0 p1 p2 p3, wound so that (p1-p0)x(p2-p0) points along n."""
        a = [p1[i] - p0[i] for i in range(3)]
        b = [p2[i] - p0[i] for i in range(3)]
        c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        pts = [p0, p1, p2, p3] if sum(c[i] * n[i] for i in range(3)) > 0 else [p3, p2, p1, p0]
        base = len(self.vertices) + 1
        self.vertices.extend(pts)
        self.faces.append((mat, [base, base + 1, base + 2, base + 3]))

    def write(self, path, materials):
        """path (.obj) and its .mtl, whose text is `materials`."""
        mtl = path[:-4] + ".mtl" if path.endswith(".obj") else path + ".mtl"
        with open(mtl, "w") as m:
            m.write(materials)
        with open(path, "w") as o:
            o.write("mtllib %s\n" % mtl.split("/")[-1])
            for v in self.vertices:
                o.write("v %g %g %g\n" % tuple(v))
            cur = None
            for mat, f in self.faces:
                if mat == "group":
                    o.write("g cell:%s\n" % f)
                    cur = None
                    continue
                if mat != cur:
                    o.write("usemtl %s\n" % mat)
                    cur = mat
                o.write("f %s\n" % " ".join(map(str, f)))
