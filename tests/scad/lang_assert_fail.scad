// A failed assert is an error with the condition's text and the message.
// expect error: assertion '(1 > 2)' failed: "too small"
assert(1 > 2, "too small");
cube(1);
