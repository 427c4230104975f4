// A name may start with digits when it is longer than the number there (OpenSCAD's
// longest-match lexer): 8bit is a name, 8 and 1e3 are numbers.
// expect echo: ECHO: 8, 8, 1000, 2.5
function 8bit() = 8;
echo(8bit(), 8, 1e3, 2.5);
