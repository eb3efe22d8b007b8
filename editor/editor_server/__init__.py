"""The parts of the field editor's server (editor/serve.py, the HTTP side and the command line)."""
