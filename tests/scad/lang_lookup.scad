// lookup() interpolates linearly and clamps at the ends.
// expect echo: ECHO: 15, 20, 10, 25
t = [[1, 10], [2, 20], [3, 30]];
echo(lookup(1.5, t), lookup(2, t), lookup(0, t), lookup(2.5, t));
