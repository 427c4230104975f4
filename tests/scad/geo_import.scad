// import() of an OFF file next to the script.
// expect volume: 1
// expect no-openscad: OpenSCAD 2021 reads OFF, but the path base differs in the compare run
import("data/unit_cube.off");
