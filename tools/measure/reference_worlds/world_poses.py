#!/usr/bin/python3
"""The poses of a Gazebo world file's models, as the world state it saves places them
(docs/worlds.md, "The authors' worlds"). Reads the file from a checkout of the authors'
repository; prints one CSV row per model: its name, the Gazebo model it is (its collision mesh's, else its materials'), and the
pose x, y, z (m), roll, pitch, yaw (rad) of the file's <state> (the model's own <pose> where the
state has none). The ground plane and Gazebo's `the_void` marker are left out.

    /usr/bin/python3 tools/measure/reference_worlds/world_poses.py \\
        CHECKOUT/monospheres/worlds/suburb3.world > worlds/suburb3/reference_poses.csv

The committed CSVs are what `Worlds.TheAuthorsWorldsPlaceEveryModelAtItsSavedPose` reads."""
import re
import sys
import xml.etree.ElementTree as ET

SKIP = {"ground_plane", "the_void"}


def model_of(model):
    """The Gazebo model a saved model is: the one whose mesh its collision uses, else the one its
    materials name (model://NAME/...)."""
    for c in model.iter("collision"):
        for u in c.iter("uri"):
            if m := re.match(r"model://([^/]+)", u.text.strip()):
                return m.group(1)
    names = {m.group(1) for u in model.iter("uri") if (m := re.match(r"model://([^/]+)", u.text.strip()))}
    return ";".join(sorted(names))


def main(path):
    world = ET.parse(path).getroot().find("world")
    state = {}
    for s in world.findall("state"):
        for m in s.findall("model"):
            state[m.get("name")] = m.find("pose").text.split()
    print("name,model,x,y,z,roll,pitch,yaw")
    for m in world.findall("model"):
        name = m.get("name")
        if name in SKIP:
            continue
        pose = state.get(name) or m.find("pose").text.split()
        print(",".join([name, model_of(m)] + pose))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: world_poses.py WORLD_FILE")
    main(sys.argv[1])
