"""meshes"""
