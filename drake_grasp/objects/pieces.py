"""Convex pieces of a user's solid for contact: CoACD's decomposition of each closed part, thin
pieces joined to a neighbour and pieces merged down to the budget, each kept to at most 64 of its
vertices and cleaned for Drake's contact; written as OBJ files and cached by the content's hash.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects import cleaning, piece_budget, repair
from drake_grasp.objects.spec import (
    COACD_THRESHOLD, CONVEXITY_TOLERANCE, MeshNote, ObjectError, _obj_text, cache_dir,
)


# Bump when loading a file gives other pieces or mass properties for the same bytes: it is part of
# the decompositions' cache key and of a mesh file's fingerprint (records are computed anew).
IMPORT_VERSION = 9  # 9: seams left open at T-junctions are split (repair.split_t_junctions)
CLEANING_VERSION = 3  # part of the cache key of decompositions: bump when cleaning changes (3: Drake's own fans)


# CoACD runs in a child process: on some meshes its C++ code aborts the whole process ("terminate
# called after throwing an instance of 'std::logic_error'": the usd-wg's chess king), which would
# end the user's command with no message. The child reads the mesh from and writes the pieces to
# .npz files; it imports only numpy and coacd.
_COACD_CHILD = """
import sys, numpy as np, coacd
data = np.load(sys.argv[1])
coacd.set_log_level("error")
result = coacd.run_coacd(coacd.Mesh(data["vertices"], data["faces"]), threshold=float(data["threshold"]),
                         max_convex_hull=int(data["max_pieces"]), preprocess_mode=str(data["preprocess"]), seed=0)
np.savez(sys.argv[2], *[np.asarray(vertices, float) for vertices, _ in result])
"""


def _coacd_in_child(mesh: trimesh.Trimesh, max_pieces: int, preprocess: str) -> list[np.ndarray] | None:
    """CoACD's convex pieces (their vertices, m) from a child process; None if the child failed."""
    with tempfile.TemporaryDirectory(prefix="coacd-") as folder:
        given, taken = Path(folder) / "mesh.npz", Path(folder) / "pieces.npz"
        np.savez(given, vertices=np.asarray(mesh.vertices, float), faces=np.asarray(mesh.faces, np.int32),
                 threshold=COACD_THRESHOLD, max_pieces=max_pieces, preprocess=preprocess)
        done = subprocess.run([sys.executable, "-c", _COACD_CHILD, str(given), str(taken)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if done.returncode != 0 or not taken.exists():
            return None
        with np.load(taken) as pieces:
            return [pieces[name] for name in sorted(pieces.files, key=lambda n: int(n.split("_")[1]))]


def _coacd_pieces(mesh: trimesh.Trimesh, max_pieces: int, label: str = "mesh") -> list[np.ndarray]:
    """CoACD's convex pieces of a closed mesh (their vertices, m): seed 0, quiet. If CoACD fails on the
    mesh as given, it is run again with its own manifold preprocessing (a remesh) on; if that fails
    too, the mesh's convex hull is its one piece for contact, with a note (mass properties come from
    the mesh itself either way)."""
    for preprocess in ("auto", "on"):
        pieces = _coacd_in_child(mesh, max_pieces, preprocess)
        if pieces:
            return pieces
    warnings.warn(f"{label}: CoACD could not decompose this part (it stopped with an error); its convex hull "
                  "is its one piece for contact", MeshNote, stacklevel=4)
    return [np.asarray(mesh.convex_hull.vertices, float)]


def _decompose(mesh: trimesh.Trimesh, key: str, max_pieces: int, label: str = "mesh") -> list[str]:
    """Convex pieces of `mesh` as OBJ files (vertices in the mesh frame), cached under `key`.

    Each piece first keeps at most `piece_budget.MAX_PIECE_VERTICES` of its vertices (a hull inside
    it, so that contact and the planner's distances stay cheap), then is cleaned for contact
    (:func:`drake_grasp.objects.cleaning.clean_pieces`: no near-duplicate vertices, no sliver
    triangles, none thinner than MIN_THICKNESS), removing at most VOLUME_TOLERANCE of the mesh's
    volume (else ObjectError). Mass properties never come from the pieces: they come from the mesh.
    """
    key = f"{key}-{piece_budget.CACHE_TAG}-c{CLEANING_VERSION}-i{IMPORT_VERSION}"
    directory = cache_dir() / "decomposed" / key
    manifest = directory / "pieces.json"
    if manifest.exists():
        names = json.loads(manifest.read_text())["pieces"]
        return [str((directory / name).resolve()) for name in names]
    hull = mesh.convex_hull
    if mesh.volume >= (1.0 - CONVEXITY_TOLERANCE) * hull.volume:
        parts = [np.asarray(hull.vertices, float)]
    else:
        warnings.warn(f"{label}: non-convex: decomposing into at most {max_pieces} convex pieces (CoACD, "
                      "seconds to minutes; cached for next time)", MeshNote, stacklevel=3)
        parts = []
        bodies = [mesh] if mesh.body_count == 1 and mesh.is_watertight else repair.closed_parts(mesh)
        # A cavity's wall (wound inward) is out of reach from outside: contact takes the outer parts.
        bodies = [body for body in bodies if body.volume > 0.0] or bodies
        for body in bodies:  # the closed parts of one object (cells, hulls): each is decomposed
            body_hull = body.convex_hull
            if body.volume >= (1.0 - CONVEXITY_TOLERANCE) * body_hull.volume:
                parts.append(np.asarray(body_hull.vertices, float))
            else:
                parts += _coacd_pieces(body, max_pieces, label)
    # Pieces too thin for contact join a neighbour, and several parts' pieces are merged down to
    # max_pieces (a merged piece is the hull of both: the added volume is bounded and said).
    parts, added = cleaning.merge_pieces(parts, max_pieces)
    if added > 0.01 * float(mesh.volume):
        warnings.warn(f"{label}: convex pieces merged to {len(parts)}: their hulls add "
                      f"{100 * added / float(mesh.volume):.1f} % to the volume for contact (not to the mass)",
                      MeshNote, stacklevel=3)
    budgeted = [piece_budget.budgeted_piece(vertices)[0] for vertices in parts]
    try:
        clean, _ = cleaning.clean_pieces(budgeted, float(mesh.volume))
    except cleaning.CleaningError as error:
        clean = _clean_shell_pieces(budgeted, float(mesh.volume), added)
        if clean is None:
            raise ObjectError(f"{label}: {error}") from None
        warnings.warn(f"{label}: a shell of thin parts ({float(mesh.volume) * 1e6:.2g} cm³ of material): "
                      f"its merged convex pieces ({sum(piece.volume for piece in clean) * 1e6:.2g} cm³) "
                      "are its solid for contact (not for the mass)", MeshNote, stacklevel=3)
    parts = [(piece.vertices, piece.faces) for piece in clean]
    # Write into a private directory, then rename it into place: a concurrent process (parallel
    # trials) either sees the complete directory or none, and the first to finish wins.
    directory.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(dir=directory.parent, prefix=key + ".tmp"))
    names = [f"piece_{index:03d}.obj" for index in range(len(parts))]
    for name, (vertices, faces) in zip(names, parts):
        (staging / name).write_text(_obj_text(vertices, faces))
    (staging / "pieces.json").write_text(json.dumps({"pieces": names}))
    try:
        os.rename(staging, directory)
    except OSError:
        shutil.rmtree(staging, ignore_errors=True)
        if not manifest.exists():
            raise
        # Another process got there first; use its pieces.
    names = json.loads(manifest.read_text())["pieces"]
    return [str((directory / name).resolve()) for name in names]


def _clean_shell_pieces(budgeted: list[np.ndarray], material_volume: float, added: float):
    """Clean pieces for a part whose plain cleaning would remove too much, or None if this does not help.

    Two things make cleaning refuse a solid that contact can still take whole:
    - a merged piece just over `cleaning.MIN_THICKNESS` can come out of the vertex budget (a hull of
      its own vertices, inside it) just under it, and would be dropped; here it joins a neighbour
      again, as `cleaning.merge_pieces` joins every thin piece;
    - a part built of thin sheets (pybullet's random_urdfs/292: 42 convex slivers 0.1-1.3 mm thick
      around a 0.9 × 6.3 × 1 cm stick, 0.29 cm³ of material) is a solid for contact only as its merged
      hulls, which hold many times the material's volume: what cleaning removes is measured against
      that solid for contact, not against the material.

    Mass properties never come from the pieces, so neither changes the mass.
    """
    pieces, volume_for_contact = budgeted, material_volume + added
    for _ in range(3):
        pieces, more = cleaning.merge_pieces(pieces, len(pieces))
        pieces = [piece_budget.budgeted_piece(vertices)[0] for vertices in pieces]
        volume_for_contact += more
        try:
            clean, _ = cleaning.clean_pieces(pieces, volume_for_contact)
        except cleaning.CleaningError:
            continue
        return clean
    return None
