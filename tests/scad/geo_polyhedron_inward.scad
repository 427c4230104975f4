// A closed shell of a polyhedron whose faces all point inward (counterclockwise seen
// from outside) is built as the volume it encloses, as OpenSCAD builds it, with a
// warning; each shell is judged alone. The wedge of legs 4 and 4 and height 2 (MCAD's
// trochoids.scad lists its wedges so) in one polyhedron with a tetrahedron listed the
// right way, united with a cube inside the wedge: 4 * 4 / 2 * 2 + 1 / 6.
// expect volume: 16.1666666666666667
// expect bbox: [0, 0, 0] [11, 4, 2]
// expect valid
// expect warning: polyhedron(): the faces of a closed shell point inward
polyhedron(points = [[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 2], [4, 0, 2], [0, 4, 2],
                     [10, 0, 0], [11, 0, 0], [10, 1, 0], [10, 0, 1]],
           faces = [[0, 2, 1], [0, 1, 3], [3, 1, 4], [3, 4, 5], [0, 3, 2], [2, 3, 5], [1, 2, 4],
                    [2, 5, 4],
                    [6, 7, 8], [6, 9, 7], [6, 8, 9], [7, 9, 8]]);
translate([1, 1, 0]) cube(1);
