"""recon3d"""
