"""windflutter.rotor"""
