# The folders of the interpreter library (mcnc_interp), relative to the repository's root: the
# top-level build and the fuzzing build (tests/fuzz) both build it from them.
set(MCNC_INTERP_FOLDERS
    channel/interp
    channel/interp/macro
    channel/interp/program
    channel/interp/parse
    channel/interp/output
    channel/interp/path
    channel/interp/cycles
    channel/interp/transform
    channel/interp/limits
    channel/interp/state)
