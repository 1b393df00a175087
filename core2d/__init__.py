"""core2d"""
