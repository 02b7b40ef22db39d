"""windflutter.mesh"""
