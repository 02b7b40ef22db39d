"""windflutter.stability"""
