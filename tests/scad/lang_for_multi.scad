// for over several variables: the first is the outer loop.
// expect echo: ECHO: 0, 0
// expect echo: ECHO: 0, 1
// expect echo: ECHO: 1, 0
// expect echo: ECHO: 1, 1
for (i = [0:1], j = [0:1]) echo(i, j);
