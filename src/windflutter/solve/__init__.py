"""windflutter.solve"""
