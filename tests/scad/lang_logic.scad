// Truth: 0, "", [] and undef are false; && and || give booleans.
// expect echo: ECHO: false, true, true, false, "b", true, false
echo(true && false, true || false, !0, !"x", 0 ? "a" : "b", [1] && 1, [] || "");
