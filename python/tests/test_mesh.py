"""Meshes from numpy arrays: the same bytes as the OBJ file of the same data
and as a trimesh-shaped object; bad arrays refused with the argument and
element named; depth and ids as arrays."""

import os
import types

import numpy as np
import pytest

import zscan

SIZE = (96, 72)
EYE = (1.2, -1.6, 1.8)


def hill(n=6):
    """A height field of (n+1)^2 vertices over [-1, 1]^2: smooth normals,
    vertex colours (floats 0..1, alpha too), texture coordinates, triangles."""
    t = np.linspace(-1.0, 1.0, n + 1)
    x, y = np.meshgrid(t, t)
    z = 0.3 * (1.0 - x * x) * (1.0 - y * y)
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    # the surface's normal: (-dz/dx, -dz/dy, 1), unit length
    dzdx, dzdy = -0.6 * x * (1.0 - y * y), -0.6 * y * (1.0 - x * x)
    normals = np.stack([-dzdx, -dzdy, np.ones_like(x)], axis=-1).reshape(-1, 3)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    colors = np.stack([(x + 1) / 2, (y + 1) / 2, 0.25 + 0 * x], axis=-1).reshape(-1, 3)
    uvs = np.stack([(x + 1) / 2, (y + 1) / 2], axis=-1).reshape(-1, 2)
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            faces.append([a, a + 1, a + n + 2])
            faces.append([a, a + n + 2, a + n + 1])
    return vertices, np.array(faces, np.int64), colors, normals, uvs


def checker():
    k = (np.arange(8)[:, None] // 2 + np.arange(8)[None, :] // 2) % 2
    tex = np.zeros((8, 8, 3), np.uint8)
    tex[k == 0] = (230, 200, 40)
    tex[k == 1] = (30, 60, 200)
    return tex


def write_obj(path, vertices, faces, colors=None, normals=None, uvs=None, texture=None,
              face_colors=None):
    """The OBJ (and MTL, PNG) of the arrays: numbers written with repr, which
    reads back as the same double."""
    d = os.path.dirname(path)
    lines = []
    if texture is not None or face_colors is not None:
        lines.append("mtllib m.mtl")
    for i, v in enumerate(vertices):
        c = "" if colors is None else " " + " ".join(repr(float(x)) for x in colors[i])
        lines.append("v " + " ".join(repr(float(x)) for x in v) + c)
    for t in uvs if uvs is not None else ():
        lines.append("vt " + " ".join(repr(float(x)) for x in t))
    for nrm in normals if normals is not None else ():
        lines.append("vn " + " ".join(repr(float(x)) for x in nrm))
    mtl = []
    if texture is not None:
        zscan.Image(texture.shape[1], texture.shape[0], texture.tobytes()).save(
            os.path.join(d, "tex.png"))
        mtl += ["newmtl textured", "Kd 1 1 1", "map_Kd tex.png"]
        lines.append("usemtl textured")
    for f, face in enumerate(faces):
        if face_colors is not None:
            mtl += ["newmtl c%d" % f, "Kd " + " ".join(repr(float(x)) for x in face_colors[f])]
            lines.append("usemtl c%d" % f)
        corner = []
        for v in face:
            v = int(v) + 1
            vt = str(v) if uvs is not None else ""
            vn = "/" + str(v) if normals is not None else ""
            corner.append(str(v) + ("/" + vt + vn if (vt or vn) else ""))
        lines.append("f " + " ".join(corner))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    if mtl:
        with open(os.path.join(d, "m.mtl"), "w") as f:
            f.write("\n".join(mtl) + "\n")


def trimesh_shaped(vertices, faces, colors, normals, uvs):
    """What trimesh.Trimesh looks like to zscan, without trimesh."""
    rgba = np.concatenate([np.floor(colors * 255 + 0.5), np.full((len(colors), 1), 255)], axis=1)
    visual = types.SimpleNamespace(kind="vertex", vertex_colors=rgba.astype(np.uint8), uv=uvs)
    return types.SimpleNamespace(vertices=vertices, faces=faces, visual=visual,
                                 vertex_normals=normals)


@pytest.mark.parametrize("shade", ["auto", "flat", "unlit", "gouraud", "phong", "normal", "id"])
def test_arrays_trimesh_and_obj_give_one_hash(tmp_path, shade):
    vertices, faces, colors, normals, uvs = hill()
    tex = checker()
    obj = str(tmp_path / "hill.obj")
    write_obj(obj, vertices, faces, colors, normals, uvs, tex)
    from_file = zscan.render(obj, size=SIZE, eye=EYE, shade=shade)
    mesh = zscan.Mesh(vertices, faces, vertex_colors=colors, normals=normals, uvs=uvs,
                      texture=tex)
    from_arrays = zscan.render(mesh, size=SIZE, eye=EYE, shade=shade)
    shaped = trimesh_shaped(vertices, faces, colors, normals, uvs)
    scene = zscan.Scene()
    scene.add(zscan.Mesh.from_trimesh(shaped, texture=tex))
    from_trimesh = scene.render(size=SIZE, eye=EYE, shade=shade)
    assert from_arrays.hash == from_file.hash == from_trimesh.hash
    # and the picture is not empty: the hill covers much of the frame
    assert from_file.stats["pixels_written"] > SIZE[0] * SIZE[1] // 4


def test_face_colours_and_polygons_equal_the_obj(tmp_path):
    vertices = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                         [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], np.float64)
    quads = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [3, 7, 6, 2], [0, 4, 7, 3], [1, 2, 6, 5]]
    colours = np.array([[0.9, 0.1, 0.1], [0.1, 0.9, 0.1], [0.1, 0.1, 0.9],
                        [0.9, 0.9, 0.1], [0.1, 0.9, 0.9], [0.5, 0.5, 0.5]])
    obj = str(tmp_path / "cube.obj")
    write_obj(obj, vertices, quads, face_colors=colours)
    for shade in ("flat", "id"):
        a = zscan.render(obj, size=SIZE, eye=(3, 2.5, 4), shade=shade)
        b = zscan.render(zscan.Mesh(vertices, quads, face_colors=colours), size=SIZE,
                         eye=(3, 2.5, 4), shade=shade)
        assert a.hash == b.hash, shade
    # a list of polygons of mixed sizes: the cube as 5 quads and 2 triangles
    mixed = quads[:5] + [[1, 2, 6], [1, 6, 5]]
    m = zscan.Mesh(vertices, mixed)
    assert zscan.render(m, size=SIZE).stats["polygons_in"] == 7


def test_objects_with_transforms_number_their_faces_in_turn():
    vertices, faces, *_ = hill(2)
    scene = zscan.Scene()
    mesh = zscan.Mesh(vertices, faces)
    left, right = np.eye(4), np.eye(4)
    left[0, 3], right[0, 3] = -1.2, 1.2
    scene.add(mesh, transform=left, name="left").add(mesh, transform=right, name="right")
    assert scene.objects == 2 and scene.faces == 2 * len(faces)
    scene.camera = {"eye": (0, -1, 5)}
    im = scene.render(size=SIZE, shade="id", depth=True)
    ids = im.ids
    assert ids.dtype == np.int32 and ids.shape == (SIZE[1], SIZE[0])
    assert ids[SIZE[1] // 2, 5] == -1  # the background between and around
    left_ids = set(ids[:, : SIZE[0] // 2].ravel()) - {-1}
    right_ids = set(ids[:, SIZE[0] // 2:].ravel()) - {-1}
    assert left_ids and max(left_ids) < len(faces) <= min(right_ids)
    assert im.depth.dtype == np.float32 and im.depth.shape == ids.shape
    assert ((im.depth < 1) == (ids >= 0)).all()
    objects = im.objects
    assert objects.dtype == np.int32 and objects.shape == ids.shape
    assert ((objects == -1) == (ids == -1)).all()
    assert (objects[ids >= len(faces)] == 1).all() and (objects[(ids >= 0) & (ids < len(faces))] == 0).all()
    assert set(np.unique(objects[:, : SIZE[0] // 2])) == {-1, 0}
    png = im._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_lights_from_python_change_the_picture():
    vertices, faces, colors, normals, uvs = hill()
    mesh = zscan.Mesh(vertices, faces, vertex_colors=colors, normals=normals)
    head = zscan.render(mesh, size=SIZE, eye=EYE, shade="phong")
    red = zscan.render(mesh, size=SIZE, eye=EYE, shade="phong",
                       lights=[zscan.Light("directional", color=(1, 0, 0), direction=(0, 0, -1))])
    assert head.hash != red.hash
    r, g, b = red.pixel(SIZE[0] // 2, SIZE[1] // 2)
    assert r > 0 and g == 0 and b == 0


V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float64)


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(vertices=np.zeros((3, 2)), faces=[[0, 1, 2]]), ValueError,
     "vertices: expected shape (N, 3), got (3, 2)"),
    (dict(vertices=[["a", "b", "c"]] * 3, faces=[[0, 1, 2]]), TypeError,
     "vertices: expected numbers, got an array of <U1"),
    (dict(vertices=np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]]), faces=[[0, 1, 2]]),
     ValueError, "vertices[1, 1]: nan is not a finite number"),
    (dict(vertices=V, faces=[[0, 1, 3]]), ValueError,
     "faces[0, 2]: vertex 3 out of range (3 vertices)"),
    (dict(vertices=V, faces=[[0, 1, 2], [0, -1, 2, 1]]), ValueError,
     "faces[1, 1]: vertex -1 out of range (3 vertices)"),
    (dict(vertices=V, faces=[[0, 1]]), ValueError,
     "faces: expected shape (M, 3), (M, 4) or (M, k), k >= 3, or a list of polygons, got shape (1, 2)"),
    (dict(vertices=V, faces=[[0, 1, 2], [0, 1]]), ValueError,
     "faces[1]: 2 corners (at least 3 needed)"),
    (dict(vertices=V, faces=np.array([[0.0, 1.0, 2.0]])), TypeError,
     "faces: expected integers, got an array of float64"),
    (dict(vertices=V, faces=[[0, 1, 2]], face_colors=[[255, 0, 300]]), ValueError,
     "face_colors[0, 2]: 300 is outside 0..255 (integers are 0..255, floats 0..1)"),
    (dict(vertices=V, faces=[[0, 1, 2]], face_colors=[[1.0, 0.5, 1.5]]), ValueError,
     "face_colors[0, 2]: 1.5 is outside 0..1 (floats are 0..1, integers 0..255)"),
    (dict(vertices=V, faces=np.array([[0, 1, 2]], np.int32), vertex_colors=np.ones((3, 3)),
          copy=False), ValueError,
     "vertex_colors: copy=False needs a C-contiguous uint8 array, got float64 (floats are "
     "converted to bytes)"),
    (dict(vertices=V, faces=[[0, 1, 2]], face_colors=[[1, 0, 0], [0, 1, 0]]), ValueError,
     "face_colors: 2 rows for 1 faces"),
    (dict(vertices=V, faces=[[0, 1, 2]], vertex_colors=np.ones((3, 5))), ValueError,
     "vertex_colors: expected shape (N, 3 or 4), got (3, 5)"),
    (dict(vertices=V, faces=[[0, 1, 2]], normals=np.array([[0, 0, 1]] * 2, np.float32)),
     ValueError, "normals: 2 rows for 3 vertices"),
    (dict(vertices=V, faces=[[0, 1, 2]], uvs=np.array([[0, 0], [1, np.inf], [0, 1]])),
     ValueError, "uvs[1, 1]: inf is not a finite number"),
    (dict(vertices=V, faces=[[0, 1, 2]], texture=np.zeros((4, 4, 3), np.uint8)), ValueError,
     "texture: needs uvs, the texture coordinates of the vertices"),
    (dict(vertices=V, faces=[[0, 1, 2]], uvs=np.zeros((3, 2)),
          texture=np.zeros((4, 4), np.uint8)), ValueError,
     "texture: expected shape (H, W, 3) or (H, W, 4), got (4, 4)"),
    (dict(vertices=V, faces=[[0, 1, 2]], uvs=np.zeros((3, 2)),
          texture=np.zeros((4, 4, 3), np.float32)), TypeError,
     "texture: expected a uint8 array, got float32"),
    (dict(vertices=np.asfortranarray(np.ones((3, 3))), faces=[[0, 1, 2]], copy=False),
     ValueError, "vertices: copy=False needs a C-contiguous float64 array, got float64 (not C-contiguous)"),
    (dict(vertices=V.astype(np.float32), faces=[[0, 1, 2]], copy=False), ValueError,
     "vertices: copy=False needs a C-contiguous float64 array, got float32"),
    (dict(vertices=V, faces=None), ValueError, "faces: a mesh needs faces, lines or points"),
    (dict(vertices=V, faces=None, lines=[[0, 3]]), ValueError,
     "lines[0, 1]: vertex 3 out of range (3 vertices)"),
])
def test_bad_arrays_name_the_argument_and_element(kwargs, error, message):
    with pytest.raises(error) as e:
        zscan.Mesh(**kwargs)
    assert str(e.value) == message


def test_arrays_in_the_librarys_layout_are_not_copied():
    faces = np.array([[0, 1, 2]], np.int32)
    m = zscan.Mesh(V, faces, copy=False)
    assert m.vertices is V
    assert np.shares_memory(m.face_vert, faces)


def test_material_colours_by_type_and_alpha_as_a_fraction():
    red = zscan.Material(color=(1.0, 0.0, 0.0), alpha=1)
    assert red.color == (255, 0, 0) and red._c.base[3] == 255
    assert zscan.Material(color=(255, 0, 0)).color == (255, 0, 0)
    assert zscan.Material(color=(1, 0, 0)).color == (1, 0, 0)  # integers are bytes
    assert zscan.Material(alpha=0.5)._c.base[3] == 128
    with pytest.raises(ValueError, match=r"^material.alpha: expected 0 .. 1, got 255$"):
        zscan.Material(alpha=255)
    with pytest.raises(ValueError, match=r"is outside 0..1"):
        zscan.Material(color=(2.0, 0.0, 0.0))


def test_bad_transforms_and_meshes_in_a_scene():
    scene = zscan.Scene()
    m = zscan.Mesh(V, [[0, 1, 2]])
    t = np.eye(4)
    t[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"^transform\[2, 1\]: nan is not a finite number$"):
        scene.add(m, transform=t)
    with pytest.raises(ValueError, match=r"^transform: expected a 4 x 4 matrix, got shape \(3, 3\)$"):
        scene.add(m, transform=np.eye(3))
    with pytest.raises(TypeError, match="^mesh: expected a zscan.Mesh or a trimesh-like mesh"):
        scene.add("cube.obj")
    assert scene.objects == 0
    scene.add(m)
    assert scene.objects == 1 and scene.faces == 1


def test_objects_of_a_file_count_what_the_command_queries(cli):
    """image.objects of a loaded scene: each object's pixels are the
    visible pixels `zscan query` prints for it."""
    import subprocess

    from conftest import CLI, CLI_ENV

    scene = zscan.load("builtin:cubes?n=2")
    objects = scene.render(size=(160, 120), shade="id").objects
    out = subprocess.run([CLI, "query", "builtin:cubes?n=2", "--size", "160x120"],
                         capture_output=True, text=True, env=CLI_ENV, check=True).stdout
    names = [line.split()[1] for line in out.splitlines() if line.startswith("object ")]
    visible = [int(line.split("visible=")[1].split()[0]) for line in out.splitlines()
               if line.startswith("object ")]
    assert len(names) == scene.objects == 8 and sum(visible) > 0
    counts = np.bincount(objects[objects >= 0].ravel(), minlength=8)
    # the command lists objects by first face, which is their order here
    assert counts.tolist() == visible
    with pytest.raises(ValueError, match=r"^Image.ids: the image was not rendered with shade='id'$"):
        scene.render(size=(16, 12)).objects


def test_normals_are_the_commands_float_for_float(tmp_path, cli):
    """image.normals is `zscan render --normals`'s PFM, bit for bit."""
    pfm = tmp_path / "n.pfm"
    r = cli("builtin:cubes?n=2", "--size", "80x60", "--normals", pfm, stats=False)
    assert r.returncode == 0, r.stderr
    data = pfm.read_bytes()
    header = b"PF\n80 60\n-1.0\n"
    assert data.startswith(header)
    theirs = np.frombuffer(data[len(header):], "<f4").reshape(60, 80, 3)[::-1]
    im = zscan.render("builtin:cubes?n=2", size=(80, 60), normals=True)
    assert im.normals.dtype == np.float32 and im.normals.shape == (60, 80, 3)
    assert im.normals.tobytes() == np.ascontiguousarray(theirs).tobytes()
    lit = np.linalg.norm(im.normals, axis=2)
    assert (lit[lit > 0] > 0.999).all() and (lit == 0).sum() > 0
    with pytest.raises(TypeError, match=r"^normals: expected True or False, got 1$"):
        zscan.render("builtin:cubes?n=2", size=(8, 6), normals=1)


def test_arrays_changed_after_the_mesh_are_named_as_arguments():
    """Arrays handed over without a copy are the caller's: a value made bad
    since is named by its argument, before the library reads it."""
    vertices = np.array(V)
    faces = np.array([[0, 1, 2]], np.int32)
    mesh = zscan.Mesh(vertices, faces, copy=False)
    faces[0, 2] = 7
    with pytest.raises(ValueError, match=r"^faces\[0, 2\]: vertex 7 out of range \(3 vertices\) "
                                         r"\(changed since the Mesh was made\)$"):
        zscan.render(mesh, size=(8, 8))
    faces[0, 2] = 2
    vertices[1, 0] = np.nan
    with pytest.raises(ValueError, match=r"^vertices\[1, 0\]: nan is not a finite number "):
        zscan.Scene().add(mesh)
    vertices[1, 0] = 1.0
    assert zscan.render(mesh, size=(8, 8)).width == 8


def test_scene_lights_and_camera_are_checked_when_set():
    scene = zscan.Scene()
    with pytest.raises(ValueError, match=r"^scene.lights: 0 lights: 1 to 16 \(None: "):
        scene.lights = []
    with pytest.raises(TypeError, match=r"^scene.lights\[1\]: expected a zscan.Light, got 'str'$"):
        scene.lights = [zscan.Light("directional", direction=(0, 0, -1)), "sun"]
    with pytest.raises(ValueError, match=r"^scene.camera: unknown key 'position' \(eye, target, "):
        scene.camera = {"position": (0, 0, 5)}
    with pytest.raises(ValueError, match=r"^scene.camera\['eye'\]: expected three numbers"):
        scene.camera = {"eye": (0, 5)}
    with pytest.raises(ValueError, match=r"^scene.camera\['fovy'\]: expected a finite number"):
        scene.camera = {"fovy": float("inf")}
    assert scene.lights is None and scene.camera == {}
    scene.camera = {"eye": [0, 0, 5], "fovy": 30}
    assert scene.camera == {"eye": (0.0, 0.0, 5.0), "fovy": 30.0}
