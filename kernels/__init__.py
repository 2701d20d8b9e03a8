"""Compiled physics of a free-standing rigid block on a moving rigid floor.

Six motion types (rest, slide, rotation, slide rotation, translation jump, rotation jump),
event-driven integration, impact laws with friction and restitution.  Importing the
package compiles nothing; the first call does (and caches on disk).
"""
from .api import (DEFAULTS, PackingError, SceneResult, record_buffer, run_cells, run_scene,
                  scene_row)

__all__ = ["DEFAULTS", "PackingError", "SceneResult", "record_buffer", "run_cells", "run_scene",
           "scene_row"]
