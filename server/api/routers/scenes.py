"""GET /api/v1/scenes: the lessons in content/, as data."""
from fastapi import APIRouter, HTTPException, Request

from ...lessons.scenes import Scene, scenes
from ..scene_urls import renamed

router = APIRouter(tags=["scenes"])


@router.get("/scenes", response_model=list[Scene], summary="All scenes (lessons) with their texts in ru, uk, en")
def list_scenes() -> list[Scene]:
    return list(scenes().values())


@router.get("/scenes/{scene_id}", response_model=Scene, summary="One scene",
            responses={301: {"description": "a former id: the scene's current address"},
                       404: {"description": "no such scene"}})
def get_scene(scene_id: str, request: Request):
    scene = scenes().get(scene_id)
    if scene is None:
        raise HTTPException(404, f"no scene '{scene_id}'")
    return renamed(request, scene_id, scene.id) or scene
