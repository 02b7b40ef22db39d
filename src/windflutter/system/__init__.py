"""The coupled turbine system: blade substructures in their rotating frames, the ground-fixed
support and drivetrain, and the multi-blade (Coleman) transformation to a time-invariant system.
"""
