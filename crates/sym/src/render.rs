//! Renders an evaluated derivation as Unicode text, LaTeX, Markdown, SymPy or JSON.
