"""Where the project's data lives, and how Drake finds it.

Models ship in ``models/`` at the top of the repository with a ``package.xml`` named ``drake_grasp``,
so they are loaded through ``package://drake_grasp/...`` URLs (never downloaded at run time).
"""

from __future__ import annotations

import pathlib

from pydrake.multibody.parsing import PackageMap, Parser

REPO_DIR = pathlib.Path(__file__).resolve().parent.parent
MODELS_DIR = REPO_DIR / "models"
DIAGRAMS_DIR = REPO_DIR / "diagrams"
PACKAGE_NAME = "drake_grasp"


def RegisterPackage(parser: Parser) -> Parser:
    """Makes ``package://drake_grasp/...`` resolve to models/ for `parser`; returns `parser`."""
    package_map: PackageMap = parser.package_map()
    if not package_map.Contains(PACKAGE_NAME):
        package_map.Add(PACKAGE_NAME, str(MODELS_DIR))
    return parser
