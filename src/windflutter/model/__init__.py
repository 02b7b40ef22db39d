"""windflutter.model"""
