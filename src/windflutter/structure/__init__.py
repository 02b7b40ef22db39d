"""windflutter.structure"""
