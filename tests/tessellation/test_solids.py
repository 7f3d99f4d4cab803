"""Voussoir solids: closed, outward-oriented, positive volume, joint faces shared exactly."""

from collections import Counter

import numpy as np
import pytest

from vaultgram.pipeline import tessellate
from vaultgram.tessellation.solids import solid_volumes


def _edges(triangles):
    return Counter((int(a), int(b)) for t in triangles for a, b in zip(t, np.roll(t, -1)))


@pytest.fixture(scope="module")
def tessellation(arch_grid):
    return tessellate(arch_grid, thickness=0.3)


def test_every_solid_is_closed_and_outward_oriented(tessellation):
    solids = tessellation.solids
    for k in range(tessellation.layout.n_voussoirs):
        count = _edges(solids.of(k))
        # closed and consistently oriented: every directed edge once, with its reverse once
        assert all(n == 1 and count.get((b, a)) == 1 for (a, b), n in count.items())
    volumes = solid_volumes(solids, tessellation.layout.n_voussoirs)
    assert (volumes > 0).all()


def test_volumes_add_up_to_the_shell(tessellation):
    """The solids tile the shell between intrados and extrados: their volumes sum to about
    thickness x mid-surface area (exactly, for a flat surface)."""
    volumes = solid_volumes(tessellation.solids, tessellation.layout.n_voussoirs)
    area = tessellation.layout.areas(tessellation.vertices).sum()
    assert volumes.sum() == pytest.approx(0.3 * area, rel=0.05)


@pytest.mark.parametrize("rows", [1, 7, 64])
def test_volumes_by_blocks_are_the_volumes_at_once(tessellation, monkeypatch, rows):
    """Triangles taken a few at a time give the volumes, bit for bit, that one block of all of them
    gives (the products and the per-solid sums are the same, in the same order)."""
    import vaultgram.tessellation.solids as module

    n = tessellation.layout.n_voussoirs
    monkeypatch.setattr(module, "VOLUME_ROWS", len(tessellation.solids.triangles))
    at_once = solid_volumes(tessellation.solids, n)
    monkeypatch.setattr(module, "VOLUME_ROWS", rows)
    assert np.array_equal(solid_volumes(tessellation.solids, n), at_once)


def test_neighbours_share_their_joint_faces_exactly(tessellation):
    solids = tessellation.solids
    owner_of = {}
    for t, k, joint in zip(solids.triangles.tolist(), solids.owner.tolist(), solids.joint.tolist()):
        if joint:
            owner_of.setdefault(frozenset(t), []).append(k)
    shared = [ks for ks in owner_of.values() if len(ks) == 2]
    alone = [ks for ks in owner_of.values() if len(ks) == 1]
    assert all(a != b for a, b in shared)
    # every joint of the layout gives two shared triangles; the rest face the boundary
    assert len(shared) == 2 * len(tessellation.layout.joints)
    assert len(alone) == 2 * int(tessellation.layout.edges.boundary.sum())


def test_flat_extrados_tops_are_planar(arch_grid):
    t = tessellate(arch_grid, thickness=0.3, flat_extrados=True)
    solids = t.solids
    n = len(t.vertices)
    for k in range(t.layout.n_voussoirs):
        tris = solids.of(k)
        tops = np.unique(tris[(tris >= 2 * n + 2 * t.layout.n_voussoirs).any(axis=1)])
        tops = tops[tops >= 2 * n + 2 * t.layout.n_voussoirs]
        p = solids.vertices[tops]
        centred = p - p.mean(axis=0)
        assert np.linalg.svd(centred, compute_uv=False)[-1] < 1e-9 * max(1.0, np.abs(p).max())
    assert (solid_volumes(solids, t.layout.n_voussoirs) > 0).all()


def test_joints_are_normal_to_the_surface(tessellation):
    tilt = tessellation.summary["joint_tilt_deg"]
    assert tilt["median"] <= 1.0 and tilt["p95"] <= 3.5
