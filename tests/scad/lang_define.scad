// -D overrides a top-level assignment (the corpus runner passes -D size=3).
// expect define: size=3
// expect echo: ECHO: 3
// expect volume: 27
size = 1;
echo(size);
cube(size);
