"""The planner's two energies, on plain arrays (docs/design.md §4.6).

Both are GraspIt!'s (src/EGPlanner/energy/contactEnergy.cpp and guidedPotentialQualityEnergy.cpp;
docs/design.md §4.6), computed from the virtual contacts of the hand (virtual_contacts.py): each
contact i has an outward unit normal n_i and a vector p_i from the contact to the closest point of
the object. GraspIt!'s constants are in millimetres: distances are converted from metres to mm at
the start of each function (``MM_PER_M``), and the energies come out in GraspIt!'s units.

* ``contact``: E = mean_i ( |p_i| + 50 (1 − n̂_i · p̂_i) ), |p| in mm ("Hand Contacts",
  CONTACT_ENERGY). Every contact counts, however far.
* ``contact-quality``: each contact gets the factor sf_i = cos(π d_i / 50 mm) + 1 when d_i ≤ 50 mm
  and n̂_i · p̂_i ≥ 0.7, else 0. When at least 3 contacts have sf > 0.25, E = −ε of the force-only
  (3-D) L1 wrench space of all contacts' friction cones scaled by their sf (friction 0.2 on palm and
  links, 1.0 on fingertips); otherwise E is the contact energy ("Contacts AND Quality",
  GUIDED_POTENTIAL_QUALITY_ENERGY). ε is 0 when the origin is not strictly inside the hull. In
  GraspIt! too, a state with 3 close contacts but no force closure scores 0 rather than its contact
  energy: the contacts scaled to 0 put the origin on the hull, and its QualEpsilon then returns 0,
  not −1 (it returns −1 only when the origin is outside).

Pure numpy (and the project's ε code in drake_grasp.quality), no Drake.
"""

from __future__ import annotations

import numpy as np

from drake_grasp.quality import friction_cone_edges, wrench_space_quality

ENERGIES = ("contact", "contact-quality")
"""Names of the energies, as the command line takes them."""

MM_PER_M = 1000.0  # GraspIt!'s lengths are in mm.

# --- docs/design.md §4.6 (contactEnergy.cpp). -----------------------------------------------------
NORMAL_WEIGHT = 50.0  # mm per unit of (1 − n̂·p̂): GraspIt!'s "d * 100.0 / 2.0".

# --- docs/design.md §4.6 (guidedPotentialQualityEnergy.cpp). --------------------------------------
QUALITY_DISTANCE_MM = 50.0  # contacts farther than this get factor 0.
QUALITY_MIN_COSINE = 0.7  # contacts whose normal is farther than ~45° from p get factor 0.
QUALITY_COUNT_FACTOR = 0.25  # a contact "counts" when its factor exceeds this,
QUALITY_MIN_CONTACTS = 3  # and the quality branch needs this many counting contacts.
QUALITY_CONE_EDGES = 8  # edges of each linearised friction cone (ε convention: docs/design.md §4.5).


def contact_energy(normals, distances, directions) -> float:
    """GraspIt!'s contact energy ("Hand Contacts").

    Args:
        normals: (N, 3) outward unit normals of the virtual contacts.
        distances: (N,) |p_i|, distance from each contact to the closest object point, m.
        directions: (N, 3) p̂_i, unit vector from each contact toward its closest object point.

    Returns:
        The mean over contacts of |p| (mm) + 50 (1 − n̂·p̂); dimension mm.
    """
    n = len(distances)
    cosine_sum = np.einsum("ij,ij->", normals, directions)
    return float(np.abs(distances).sum() * MM_PER_M + NORMAL_WEIGHT * (n - cosine_sum)) / n


def contact_energy_from_points(points, normals, closest_points) -> float:
    """:func:`contact_energy` from contact points and the object's closest points (m).

    p = closest − point. A contact that touches the object (p = 0) has no direction and counts
    with n̂·p̂ = 0 here; the planner calls :func:`contact_energy` with the object's surface normal
    as the direction instead, which is the limit of p̂ as the contact approaches the surface.
    """
    p = np.asarray(closest_points, dtype=float) - np.asarray(points, dtype=float)
    length = np.linalg.norm(p, axis=1)
    directions = np.divide(p, length[:, None], out=np.zeros_like(p), where=length[:, None] > 0.0)
    return contact_energy(np.asarray(normals, dtype=float), length, directions)


def quality_scale(distances, cosines) -> np.ndarray:
    """GraspIt!'s potential-quality factor of each contact.

    Args:
        distances: (N,) contact-to-object distances, m.
        cosines: (N,) n̂·p̂ of each contact.

    Returns:
        (N,) sf = cos(π d / 50 mm) + 1 where d ≤ 50 mm and n̂·p̂ ≥ 0.7, else 0 (in [0, 2]).
    """
    d_mm = np.abs(np.asarray(distances, dtype=float)) * MM_PER_M
    cosines = np.asarray(cosines, dtype=float)
    sf = np.cos(np.pi * d_mm / QUALITY_DISTANCE_MM) + 1.0
    return np.where((d_mm <= QUALITY_DISTANCE_MM) & (cosines >= QUALITY_MIN_COSINE), sf, 0.0)


def force_space_epsilon(edges, scale) -> float:
    """ε of the force-only (3-D) L1 wrench space of scaled friction cones.

    Args:
        edges: (N, m, 3) friction-cone edges of the contacts (normal component 1), in any frame
            (ε does not depend on it), e.g. from ``drake_grasp.quality.friction_cone_edges``.
        scale: (N,) factors the cones are scaled by; contacts with factor 0 add nothing.

    Returns:
        Distance from the origin to the nearest facet of the hull of all scaled cone edges, or 0
        when the origin is not strictly inside (or the edges span less than 3-D).
    """
    scale = np.asarray(scale, dtype=float)
    used = scale > 0.0
    if np.count_nonzero(used) == 0:
        return 0.0
    edges = np.asarray(edges, dtype=float)[used]
    forces = (edges * scale[used][:, None, None]).reshape(-1, 3)
    # Cheap rejection: when every force has a non-negative component along some direction (the
    # mean force, or a contact's cone axis), the origin is not strictly inside the hull.
    directions = np.vstack((forces.mean(axis=0), edges.mean(axis=1)))
    if np.any(np.all(forces @ directions.T >= 0.0, axis=0)):
        return 0.0
    return wrench_space_quality(forces).epsilon


def contact_quality_energy(normals, distances, directions, friction, cone_edges=None) -> float:
    """GraspIt!'s "Contacts AND Quality" energy.

    Args:
        normals: (N, 3) outward unit normals of the virtual contacts.
        distances: (N,) contact-to-object distances, m.
        directions: (N, 3) unit vectors from each contact toward its closest object point.
        friction: (N,) friction coefficient of each contact.
        cone_edges: (N, m, 3) the contacts' friction-cone edges, in any frame, or a function
            returning them (called only when needed); default: built from ``normals`` and
            ``friction`` with ``QUALITY_CONE_EDGES`` edges. GraspIt!'s virtual
            contacts carry their edges in their link frames; the planner passes edges built in the
            hand frame, so the linearised cones turn with the hand.

    Returns:
        −ε (≤ 0) of the sf-scaled force space when at least 3 contacts have sf > 0.25, else the
        contact energy (> 0).
    """
    cosines = np.einsum("ij,ij->i", normals, directions)
    sf = quality_scale(distances, cosines)
    if np.count_nonzero(sf > QUALITY_COUNT_FACTOR) < QUALITY_MIN_CONTACTS:
        n = len(cosines)
        return float(np.abs(distances).sum() * MM_PER_M + NORMAL_WEIGHT * (n - cosines.sum())) / n
    if callable(cone_edges):
        cone_edges = cone_edges()
    elif cone_edges is None:
        cone_edges = friction_cone_edges(np.asarray(normals, dtype=float), np.asarray(friction, dtype=float),
                                         QUALITY_CONE_EDGES)
    return -force_space_epsilon(cone_edges, sf)
