"""The assembler's passes, one module each."""
