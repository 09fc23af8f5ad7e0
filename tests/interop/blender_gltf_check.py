"""Runs inside Blender (blender --background --factory-startup --python THIS -- ARGS).

Imports a glTF file with Blender's own importer, steps the scene to each sample's frame
(subframes included), and writes the world positions of the animated mesh's vertices.

Usage: blender ... --python blender_gltf_check.py -- FILE.glb SAMPLES.json RESULT.json
SAMPLES.json: {"frames": [f, ...]}; RESULT.json: {"fps": ..., "positions": [[[x,y,z],...],...]}
"""
import json
import sys

import bpy


def main():
    glb, samples_path, result_path = sys.argv[sys.argv.index("--") + 1:][:3]
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    # Shading "FLAT": Debian 12's Blender 3.4 importer, with its default "NORMALS", calls
    # numpy.bool, which Debian's numpy 1.24 no longer has, and fails on every mesh.
    bpy.ops.import_scene.gltf(filepath=glb, import_shading="FLAT")
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        raise SystemExit("expected one mesh object, found %d" % len(meshes))
    body = meshes[0]
    scene = bpy.context.scene
    fps = scene.render.fps / scene.render.fps_base
    with open(samples_path) as f:
        frames = json.load(f)["frames"]
    positions = []
    for frame in frames:
        whole = int(frame // 1)
        scene.frame_set(whole, subframe=frame - whole)
        world = body.matrix_world.copy()
        positions.append([list(world @ v.co) for v in body.data.vertices])
    action = body.animation_data.action if body.animation_data else None
    with open(result_path, "w") as f:
        json.dump({"fps": fps, "positions": positions,
                   "action": action.name if action else None,
                   "frame_range": list(action.frame_range) if action else None}, f)


main()
