// A closed polyhedron whose faces all point inward (counterclockwise seen from
// outside) is built as the volume it encloses, as OpenSCAD builds it, with a warning:
// the wedge of legs 4 and 4 and height 2 (MCAD's trochoids.scad lists its wedges so),
// united with a cube inside it: 4 * 4 / 2 * 2 = 16.
// expect volume: 16
// expect bbox: [0, 0, 0] [4, 4, 2]
// expect valid
// expect warning: polyhedron(): the faces point inward
polyhedron(points = [[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 2], [4, 0, 2], [0, 4, 2]],
           faces = [[0, 2, 1], [0, 1, 3], [3, 1, 4], [3, 4, 5], [0, 3, 2], [2, 3, 5], [1, 2, 4],
                    [2, 5, 4]]);
translate([1, 1, 0]) cube(1);
