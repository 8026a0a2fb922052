# Manual check that Blender opens mocapdb's BVH export and poses it as mocapdb's FK does.
# Not part of the test suite (Blender is not a project dependency). Usage:
#   apt-get install blender
#   build/release/tools/mocapdb convert ../shared/datasets/cmu-asfamc/16_15.amc -o /tmp/bl/16_15.bvh
#   blender -b --python scripts/blender_import_check.py
# Prints the bone count, frame range and three joints' world positions at frames 1, 200 and 471;
# Blender's Z-up (x, y, z) equals mocapdb's Y-up (x, -z, y); compare with `mocapdb` FK positions.
import bpy, sys, builtins
# Debian's Blender 3.4 BVH importer opens files with mode 'rU', which Python 3.11 refuses (the same
# for any BVH file); strip the obsolete 'U' so the importer itself runs unchanged.
_open = builtins.open
builtins.open = lambda f, mode='r', *a, **k: _open(f, mode.replace('U', ''), *a, **k)
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_anim.bvh(filepath="/tmp/bl/16_15.bvh", global_scale=1.0, frame_start=1, use_fps_scale=False, rotate_mode='NATIVE', axis_forward='-Z', axis_up='Y')
arm = [o for o in bpy.context.scene.objects if o.type == 'ARMATURE'][0]
print("BONES", len(arm.data.bones))
act = arm.animation_data.action
print("FRAMES", act.frame_range[0], act.frame_range[1])
scene = bpy.context.scene
for f in (1, 200, 471):
    scene.frame_set(f)
    for name in ("lhand", "rtoes", "head"):
        pb = arm.pose.bones[name]
        p = arm.matrix_world @ pb.head
        print("POS", f, name, p.x, p.y, p.z)
