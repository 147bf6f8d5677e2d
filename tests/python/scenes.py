"""Scenes the tests derive from data/: written once per session into a temporary folder."""
import os
import tempfile


def three_disk_in_rad_s(path):
    """data/three_disk_rotor.toml with its [speeds] in rad/s (0 to 15000 rpm written as rad/s): for tests whose
    speeds are written in rad/s, the unit a call takes by default for such a scene (its [speeds] units)."""
    text = open(path).read()
    rad = text.replace('to = 15000\ncount = 151\nunits = "rpm"', 'to = 1570.796\ncount = 151\nunits = "rad/s"')
    assert rad != text, "data/three_disk_rotor.toml: its [speeds] are no longer 0 to 15000 rpm in 151 speeds"
    out = os.path.join(tempfile.mkdtemp(), "three_disk_rotor_rad_s.toml")
    with open(out, "w") as f:
        f.write(rad)
    return out
