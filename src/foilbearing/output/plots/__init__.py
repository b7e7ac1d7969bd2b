"""Figures. Imported lazily: physics modules never import matplotlib; each function returns its Figure."""
