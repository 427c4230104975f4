// .x .y .z on vectors; an index past the end is undef.
// expect echo: ECHO: 1, 2, 3, undef
v = [1, 2, 3];
echo(v.x, v.y, v.z, v[5]);
