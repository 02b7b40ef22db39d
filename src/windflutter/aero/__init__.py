"""windflutter.aero"""
