"""zscan.Device, a culling experiment's tools: draws equal to render()'s,
occlusion queries with the modelled latency, the clock and the counters."""

import numpy as np
import pytest

import zscan

SIZE = (64, 48)
WALL = zscan.Mesh(np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float),
                  [[0, 1, 2, 3]], face_colors=[[200, 100, 50]])


def frame(latency_ns=20000.0, boxes=()):
    dev = zscan.Device(SIZE, clock={"query_latency_ns": latency_ns})  # render's background
    dev.camera(eye=(0, 0, 8), target=(0, 0, 0), up=(0, 1, 0), fovy=45, near=0.1, far=1000)
    dev.clear()
    dev.draw(WALL)
    queries = [dev.query_box(lo, hi) for lo, hi in boxes]
    return dev, queries


def test_a_draw_is_what_render_draws():
    dev, _ = frame()
    im = dev.finish()
    ref = zscan.render(WALL, size=SIZE, eye=(0, 0, 8), target=(0, 0, 0), up=(0, 1, 0), fovy=45,
                       near=0.1, far=1000)
    assert ref.pixel(0, 0) == (0x1E, 0x22, 0x28) and zscan.RENDER_BACKGROUND == 0x1E2228
    assert im.hash == ref.hash
    assert dev.stats == ref.stats
    ids = dev.id_buffer
    assert ids.dtype == np.uint32 and ids.shape == (SIZE[1], SIZE[0])
    assert ids[24, 32] == 0 and ids[0, 0] == 0xFFFFFFFF
    assert dev.depth_buffer[0, 0] == 0xFFFFFFFF and dev.depth_buffer[24, 32] < 0xFFFFFFFF
    assert int((ids == 0).sum()) == dev.stats["pixels_written"]


def test_queries_count_what_the_wall_leaves_and_wait_for_the_latency():
    hidden, beside = ((-1, -1, -5), (1, 1, -3)), ((3, -1, -1), (4, 1, 1))
    dev, (qh, qv) = frame(boxes=(hidden, beside))
    assert dev.query_ready(qh) is False  # 20 us have not passed on the modelled CPU
    assert dev.query_result(qh) == 0
    assert dev.clock["stalls"] == 1 and dev.clock["stall_ps"] > 0
    # qv ended after qh on the GPU: its answer comes later still
    assert dev.query_ready(qv) is False
    samples = dev.query_result(qv)
    assert samples > 0 and dev.clock["stalls"] == 2 and dev.clock["query_waits"] == 2
    # the same frame again: the same samples and the same modelled time
    again, (_, qv2) = frame(boxes=(hidden, beside))
    assert again.query_result(qv2) == samples
    again.query_result(_)
    assert again.frame_ps == dev.frame_ps > 0

    # no latency, no stall: a wait is for the queued GPU work alone (sync)
    quick, (qh0, qv0) = frame(latency_ns=0, boxes=(hidden, beside))
    assert quick.query_result(qh0) == 0 and quick.query_result(qv0) == samples
    assert quick.clock["stalls"] == 0 and quick.clock["stall_ps"] == 0
    assert quick.frame_ps < dev.frame_ps
    # CPU work reported moves the CPU clock
    before = quick.clock["cpu_ps"]
    quick.cpu_work("node", 1000)
    assert quick.clock["cpu_ps"] > before


def test_a_query_not_begun_is_refused():
    dev, (q,) = frame(boxes=(((3, -1, -1), (4, 1, 1)),))
    with pytest.raises(ValueError, match=r"^q: query 1 was not begun in this frame \(0 .. 0 were\)$"):
        dev.query_result(1)
    dev.clear()
    with pytest.raises(ValueError, match=r"^q: query 0 was not begun in this frame \(none was\)$"):
        dev.query_ready(q)


def test_normals_and_ids_from_the_device():
    hill = zscan.Mesh(np.array([[-2, -2, 0], [2, -2, 0], [0, 2, 1]], float), [[0, 1, 2]],
                      normals=[[0, 0, 1], [0, 0, 1], [0, 0, 1]])
    dev = zscan.Device(SIZE, normals=True)  # normals need a shading of attributes
    dev.camera(eye=(0, 0, 8))
    dev.clear()
    dev.draw(hill, id_base=41)
    im = dev.finish()
    assert set(np.unique(dev.id_buffer)) == {41, 0xFFFFFFFF}
    assert im.normals.shape == (SIZE[1], SIZE[0], 3) and im.normals.dtype == np.float32
    inside = dev.id_buffer == 41
    assert (np.linalg.norm(im.normals[inside], axis=1) > 0.999).all()
    assert (im.normals[~inside] == 0).all()
    ids = zscan.Device(SIZE, shade="id")
    ids.camera(eye=(0, 0, 8))
    ids.clear()
    ids.draw(hill, id_base=41)
    im = ids.finish()
    assert set(np.unique(im.ids)) == {-1, 41}
    with pytest.raises(ValueError, match=r"^Image.objects: only a Scene's render knows"):
        im.objects
    assert zscan.Device(SIZE).finish().normals is None


def test_bad_device_arguments():
    with pytest.raises(ValueError, match=r"^size: 0x48: each side must be 1 to 16384$"):
        zscan.Device((0, 48))
    with pytest.raises(ValueError, match=r"^algo: expected 'zbuffer', 'scanline', got 'depthsort'$"):
        zscan.Device(SIZE, algo="depthsort")
    with pytest.raises(ValueError, match=r"^clock: unknown parameter 'latency'"):
        zscan.Device(SIZE, clock={"latency": 1})
    dev = zscan.Device(SIZE)
    with pytest.raises(zscan.Error, match="eye and target coincide"):
        dev.camera(eye=(0, 0, 0), target=(0, 0, 0))
    with pytest.raises(TypeError, match=r"^mesh: expected a zscan.Mesh, got 'str'$"):
        dev.draw("wall.obj")
    with pytest.raises(ValueError, match=r"^transform\[0, 3\]: inf is not a finite number$"):
        t = np.eye(4)
        t[0, 3] = np.inf
        dev.draw(WALL, transform=t)
    scan = zscan.Device(SIZE, algo="scanline")
    with pytest.raises(ValueError, match="scanline mode keeps no full-frame buffers"):
        scan.depth_buffer
