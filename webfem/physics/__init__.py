"""Closed-form physics of the paper: Eq. 21 gap, asperity contact, friction. No meshes here."""
