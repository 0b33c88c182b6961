from enum import StrEnum

class ConfigurationShoulder(StrEnum):
    BACK = "back"
    FRONT = "front"

    def __str__(self) -> str:
        return str(self.value)
