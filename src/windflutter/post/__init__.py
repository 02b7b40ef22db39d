"""windflutter.post"""
