// A module's assignments are its own; the file's variable is unchanged.
// expect echo: ECHO: 2
// expect echo: ECHO: 1
x = 1;
module m() { x = 2; echo(x); }
m();
echo(x);
