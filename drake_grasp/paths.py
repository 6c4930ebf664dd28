"""Where the project's data lives, and how Drake finds it.

The hand, arm and table models live in ``models/`` at the top of the repository (with a
``package.xml`` named ``drake_grasp``) and the scenario files in ``diagrams/``. The package reaches
both through ``drake_grasp/models`` and ``drake_grasp/diagrams``, links to those folders, so that the
same paths work in a source checkout, an editable install and an installed wheel (the wheel carries
the folders' files as package data, see pyproject.toml). Models are loaded through
``package://drake_grasp/...`` URLs and never downloaded at run time.
"""

from __future__ import annotations

import pathlib

from pydrake.multibody.parsing import PackageMap, Parser

PACKAGE_DIR = pathlib.Path(__file__).resolve().parent
MODELS_DIR = pathlib.Path(__file__).parent / "models"
DIAGRAMS_DIR = pathlib.Path(__file__).parent / "diagrams"
PACKAGE_NAME = "drake_grasp"


def RegisterPackage(parser: Parser) -> Parser:
    """Makes ``package://drake_grasp/...`` resolve to models/ for `parser`; returns `parser`."""
    package_map: PackageMap = parser.package_map()
    if not package_map.Contains(PACKAGE_NAME):
        package_map.Add(PACKAGE_NAME, str(MODELS_DIR.resolve()))
    return parser
