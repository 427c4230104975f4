// String escapes: tab, \x, \u.
// expect echo: ECHO: "a	b", "A", "☺"
echo("a\tb", "\x41", "\u263A");
