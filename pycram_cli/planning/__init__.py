"""Motion planning: how the robot reaches, moves, grasps, places, opens drawers and looks, every motion
collision-checked, without carrying anything out.

The floor between `reasoning/` (what holds in the world: IK, visibility, stability) and the executors
that act (`process_modules/`); `locations/` and `designators/` ask it what would work. By job:

* `motion.py`     collision-checked motions of joints along a straight joint-space path
* `paths.py`      ways around what is in the way (via poses, named poses, a joint-space search)
* `reach.py`      the tool to a pose (inverse kinematics near the arm's configuration, straight moves), rest poses,
                  gripper values
* `grasps.py`     grasps from the object's own frame
* `pick_place.py` the grasp and the place an arm can carry out, and the object settling
* `drawers.py`    grasping a drawer handle and following it
* `head.py`       pointing the camera, however it is mounted
* `contacts.py`   what the robot penetrates right now (what it stands on is support)
"""
