"""Where the workbench's resources are (icons, task panel .ui files, translations)."""

import os

REPO_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESOURCES_DIR = os.path.join(REPO_DIR, "resources")
ICON_DIR = os.path.join(RESOURCES_DIR, "icons")
UI_DIR = os.path.join(RESOURCES_DIR, "ui")
TRANSLATIONS_DIR = os.path.join(RESOURCES_DIR, "translations")
MACHINES_DIR = os.path.join(RESOURCES_DIR, "machines")


def icon(name: str) -> str:
    """Path of ``resources/icons/<name>.svg``."""
    return os.path.join(ICON_DIR, name + ".svg")


def ui(name: str) -> str:
    """Path of ``resources/ui/<name>.ui``."""
    return os.path.join(UI_DIR, name + ".ui")
